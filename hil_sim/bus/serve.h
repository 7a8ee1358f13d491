/* `hil_sim serve`: the device firmware (fs_app on the host port's simulator CAN backend) against
 * the simulated plant in real time (times a speed factor), with the CAN bus served to clients on
 * 127.0.0.1 over the socketcand protocol (scand.h) through the bus timing model (bus_model.h). */
#ifndef SERVE_H
#define SERVE_H

/** Entry point of the subcommand (argv without "hil_sim serve"); returns the exit status. */
int bus_cmd_serve(int argc, char **argv);

#endif /* SERVE_H */
