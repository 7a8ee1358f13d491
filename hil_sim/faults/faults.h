/* `hil_sim faults`: every fault scenario of hil_sim/scenarios/faults (one .toml file each) injected into the
 * full device application in lockstep (fault_rig.h); writes the table of docs/safety.md
 * (detection time, time to zero force, worst force, latched, lost, pass) as markdown and JSON.
 * Exit status 0 when every row passes, 1 otherwise, 2 on a usage/scenario error. */
#ifndef FAULTS_H
#define FAULTS_H

/** Entry point of the subcommand (argv without "hil_sim faults"). */
int faults_cmd(int argc, char **argv);

#endif /* FAULTS_H */
