/* The processor-in-the-loop image of the MPS2 boards (fs_pil.elf, started by `hil_sim pil`):
 * the port's main loop (cm_main, firmware/ports/mps2) over the simulator's plant (pil_plant.c). */
#include "pil_plant.h"

int main(void)
{
    return cm_main(&pil_plant);
}
