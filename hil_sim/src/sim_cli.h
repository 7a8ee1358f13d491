/* hil_sim subcommands. Each takes (argc, argv) after the subcommand name and returns the exit
 * status: 0 ok, 1 run-time failure, 2 bad usage or bad input file. */
#ifndef SIM_CLI_H
#define SIM_CLI_H

/** `hil_sim run SCENARIO [options]`: run one scenario, write the CSV log and JSON summary. */
int sim_cmd_run(int argc, char **argv);

#endif /* SIM_CLI_H */
