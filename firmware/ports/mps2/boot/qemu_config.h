/* boot_config_t of the qemu demo (layout in qemu_layout.h), shared by bootloader and app. */
#ifndef QEMU_CONFIG_H
#define QEMU_CONFIG_H

#include "boot.h"

/** Build the flash devices, attach the state record store, fill *cfg. Returns the nvm status. */
int ql_config(boot_config_t *cfg);

/** Printable name of a status code (for the console). */
const char *ql_status_name(boot_status_t st);

#endif /* QEMU_CONFIG_H */
