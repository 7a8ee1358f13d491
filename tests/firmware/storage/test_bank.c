/* Skill bank: a stored skill is validated into the inactive buffer and swapped in only at a
 * tick boundary while idle; a rejected or unreadable skill leaves the active one untouched. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fls_ram.h"
#include "vectors_io.h"
#include "nvm_bank.h"

#define SECTOR 8192u
static uint8_t g_mem[SECTOR * 8u];
static uint8_t g_scratch[SECTOR];

static void test_swap_at_idle_tick_only(void **state)
{
    (void)state;
    fls_ram_t ram;
    fls_dev_t dev;
    fls_ram_init(&ram, &dev, g_mem, SECTOR, 8, 4);
    nvm_t n;
    assert_int_equal(nvm_init(&n, &dev), NVM_OK);
    static uint8_t a[SECTOR], b[SECTOR];
    const uint32_t la = tv_read("press_n10_lwr_hold.skill", a, sizeof a);
    assert_true(la > 0u && la < sizeof a);
    const uint32_t lb = tv_read("engrave_n50_ridge_release.skill", b, sizeof b);
    assert_true(lb > 0u && lb < sizeof b);
    assert_int_equal(nvm_write(&n, 0, a, la), NVM_OK);
    assert_int_equal(nvm_write(&n, 1, b, lb), NVM_OK);

    nvm_bank_t *bank = malloc(sizeof *bank);   /* test only: ~100 KB in double */
    assert_non_null(bank);
    nvm_bank_init(bank);
    assert_null(nvm_bank_active(bank));
    assert_false(nvm_bank_tick(bank, true));

    fs_status_t ps;
    assert_int_equal(nvm_bank_stage(bank, &n, 0, g_scratch, sizeof g_scratch, &ps), NVM_OK);
    assert_int_equal(ps, FS_OK);
    assert_null(nvm_bank_active(bank));           /* not before the tick */
    assert_false(nvm_bank_tick(bank, false));     /* not while executing */
    assert_null(nvm_bank_active(bank));
    assert_true(nvm_bank_tick(bank, true));
    const skill_t *s0 = nvm_bank_active(bank);
    assert_non_null(s0);
    assert_int_equal(s0->dmp.n_kernels, 10);
    assert_int_equal(bank->active_slot, 0);

    /* stage slot 1 while slot 0 runs: the active skill is unchanged until an idle tick */
    assert_int_equal(nvm_bank_stage(bank, &n, 1, g_scratch, sizeof g_scratch, &ps), NVM_OK);
    assert_ptr_equal(nvm_bank_active(bank), s0);
    assert_int_equal(nvm_bank_active(bank)->dmp.n_kernels, 10);
    assert_false(nvm_bank_tick(bank, false));
    assert_true(nvm_bank_tick(bank, true));
    assert_int_equal(nvm_bank_active(bank)->dmp.n_kernels, 50);
    assert_int_equal(nvm_bank_active(bank)->end_policy, SKILL_END_RELEASE);
    assert_int_equal(bank->active_slot, 1);

    /* a stored image that fails skill_parse (valid record, bad skill CRC) is refused */
    b[200] ^= 0x01u;
    assert_int_equal(nvm_write(&n, 2, b, lb), NVM_OK);
    assert_int_equal(nvm_bank_stage(bank, &n, 2, g_scratch, sizeof g_scratch, &ps), NVM_ERR_PAYLOAD);
    assert_int_equal(ps, FS_ERR_SKILL_CRC);
    assert_false(nvm_bank_tick(bank, true));
    assert_int_equal(nvm_bank_active(bank)->dmp.n_kernels, 50);
    /* empty slot, too small a scratch buffer */
    assert_int_equal(nvm_bank_stage(bank, &n, 3, g_scratch, sizeof g_scratch, &ps), NVM_ERR_EMPTY);
    assert_int_equal(nvm_bank_stage(bank, &n, 0, g_scratch, 100, &ps), NVM_ERR_BUFFER);
    assert_false(nvm_bank_tick(bank, true));
    assert_int_equal(bank->active_slot, 1);
    free(bank);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_swap_at_idle_tick_only),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
