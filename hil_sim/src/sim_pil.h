/* `hil_sim pil`: the processor-in-the-loop device, the product's Cortex-M image under qemu with
 * its UART on a local TCP port (SLCAN: python-can's slcan interface, socket://127.0.0.1:P). */
#ifndef SIM_PIL_H
#define SIM_PIL_H

/** Entry of the subcommand (argv after "pil"); exit status. */
int sim_cmd_pil(int argc, char **argv);

#endif /* SIM_PIL_H */
