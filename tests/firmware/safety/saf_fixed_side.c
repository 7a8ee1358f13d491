/* fs_safety_fx behind saf_fixed_side.h. */
#include "saf_fixed_side.h"

#include <string.h>

#include "saf.h"

static saf_config_t cfg;
static saf_state_t st;

void side_fx_reset(const side_cfg_t *c)
{
    saf_default_config(&cfg);
    for (unsigned a = 0; a < SAF_AXES; a++) {
        cfg.lim.axis[a].force_max_N = (fs_real_t)c->force_max_N;
        cfg.lim.axis[a].slew_max_N = (fs_real_t)c->slew_max_N;
        cfg.lim.axis[a].contact_force_max_N = (fs_real_t)c->contact_force_max_N;
        cfg.sen.axis[a].spike_N = (fs_real_t)c->spike_N;
        cfg.sen.axis[a].jump_m = (fs_real_t)c->jump_m;
        cfg.sen.axis[a].stuck_ticks = c->stuck_ticks;
    }
    cfg.lim.slew_fault_ticks = c->slew_fault_ticks;
    cfg.wdg.timeout_ms = c->timeout_ms;
    saf_init(&st);
    saf_prepare(&cfg, &st);
}

void side_fx_step(const side_in_t *in, side_out_t *out)
{
    out->clear_result = 0u;
    if (in->clear) {
        out->clear_result = (uint16_t)saf_clear_request(&cfg, &st, in->now_ms);
    }
    saf_input_t s;
    memset(&s, 0, sizeof s);
    s.tick = in->tick;
    s.now_ms = in->now_ms;
    s.host_frame = in->host_frame;
    for (unsigned a = 0; a < SAF_AXES; a++) {
        s.meas[a].pos_m = in->pos_q24[a];
        s.meas[a].vel_mps = in->vel_q24[a];
        s.meas[a].force_N = in->force_q16[a];
        s.force_req_N[a] = in->req_q16[a];
    }
    saf_output_t o;
    saf_step(&cfg, &st, &s, &o);
    for (unsigned a = 0; a < SAF_AXES; a++) {
        out->cmd_q16[a] = o.force_cmd_N[a];
    }
    out->enable = o.actuator_enable;
    out->stopping = o.stopping;
    out->fault_code = o.fault_code;
    out->cause_mask = o.cause_mask;
    out->lim_flags = o.lim_flags;
}
