/* ct_timestep.h -- part of contact.h (to be filled by its concept). */
#ifndef CT_TIMESTEP_H
#define CT_TIMESTEP_H
#endif
