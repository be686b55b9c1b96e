/* ct_force.h -- part of contact.h (to be filled by its concept). */
#ifndef CT_FORCE_H
#define CT_FORCE_H
#endif
