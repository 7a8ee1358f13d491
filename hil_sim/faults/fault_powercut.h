/* `hil_sim powercut`: on the lockstep rig (fault_rig.h, the full device on the host port), one run
 * per flash erase/program of (a) a skill download into slot 1 over UDS, (b) a firmware update
 * (level 3, RequestDownload of the image into the inactive slot, mark-test, ECUReset, the test
 * boot's self-test and confirmation) and (c) the third wrong key at level 1 after two (the
 * wrong-key record's write of the lockout): the power is cut just after operation i (every later
 * operation fails, changing nothing: hal_host_flash_cut_after), then comes back and the device
 * boots. Checked each time: the old or the new skill / firmware, complete (CRC and parse; hash and
 * tag), the other slot and the regions not written untouched (hashes), the boot state confirmed
 * with at most one test boot, the SecurityAccess record (wrong-key counter) as it was; for (c)
 * the record holds the two wrong keys or the lockout, never fewer, and the device's seed answer
 * after the power-up delay follows it. Prints the
 * count of cut points and the outcome table (docs/safety.md); exit 1 on any bad outcome. */
#ifndef FAULT_POWERCUT_H
#define FAULT_POWERCUT_H

/** Entry point of the subcommand (argv without "hil_sim powercut"). */
int powercut_cmd(int argc, char **argv);

#endif /* FAULT_POWERCUT_H */
