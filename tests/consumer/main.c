/* A program outside the tree that uses the installed firmware libraries: parse a skill image
 * (forceskill::core), convert it to fixed point (forceskill::fixed), protect and check a CAN
 * frame (forceskill::proto), with the codes and identifiers of forceskill::base.
 * usage: consumer SKILL_FILE   prints one line and exits 0 when every step agrees */
#include <stdio.h>
#include <string.h>

#include "dmpfx.h"
#include "e2e.h"
#include "fs_status.h"
#include "proto_ids.h"
#include "skill.h"

static uint8_t image[SKILL_IMAGE_MAX];

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: consumer SKILL_FILE\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (f == NULL) {
        fprintf(stderr, "consumer: cannot open %s\n", argv[1]);
        return 2;
    }
    const size_t n = fread(image, 1u, sizeof(image), f);
    (void)fclose(f);

    static skill_t skill;
    const fs_status_t parsed = skill_parse(image, (uint32_t)n, &skill);
    image[n - 1u] ^= 0x01u; /* one flipped bit: the CRC must catch it */
    static skill_t bad;
    const fs_status_t corrupted = skill_parse(image, (uint32_t)n, &bad);

    static dmpfx_model_t fx;
    const fs_status_t converted = dmpfx_from_model(&skill.dmp, &fx);

    can_frame_t frame;
    memset(&frame, 0, sizeof(frame));
    frame.id = PROTO_ID_STATUS(3u);
    frame.len = 8u;
    e2e_protect(&frame, 5u);
    e2e_rx_t rx;
    e2e_rx_reset(&rx);
    const proto_status_t first = e2e_check(&rx, &frame);
    const proto_status_t replay = e2e_check(&rx, &frame);

    const int ok = parsed == FS_OK && corrupted == FS_ERR_SKILL_CRC && converted == FS_OK &&
                   frame.id == 0x183u && first == PROTO_OK && replay == PROTO_ERR_E2E_COUNTER;
    printf("consumer: kernels=%u parse=%d corrupted=%d fixed=%d status_id=0x%03X e2e=%d,%d %s\n",
           (unsigned)skill.dmp.n_kernels, (int)parsed, (int)corrupted, (int)converted,
           (unsigned)frame.id, (int)first, (int)replay, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
