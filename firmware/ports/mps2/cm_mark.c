/* Count markers of the Cortex-M images (cm_port.h): empty, never inlined. */
#include "cm_port.h"

void cm_port_mark_begin(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_end(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_idle(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_execute(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_upload(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_other(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_teach(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_fwupdate(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_port_mark_fault(void)
{
    __asm__ volatile("" ::: "memory");
}
