/* The processor-in-the-loop plant of the MPS2 images: the simulator's plant behind the
 * interface the port declares for its main loop (firmware/ports/mps2/cm_plant.h). */
#ifndef PIL_PLANT_H
#define PIL_PLANT_H

#include "cm_plant.h"

/** The plant of `hil_sim pil`'s image (pil_plant.c), for cm_main. */
extern const cm_plant_t pil_plant;

#endif /* PIL_PLANT_H */
