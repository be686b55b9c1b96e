/* ct_friction.h -- part of contact.h (to be filled by its concept). */
#ifndef CT_FRICTION_H
#define CT_FRICTION_H
#endif
