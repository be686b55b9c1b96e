/* ct_narrow.h -- part of contact.h (to be filled by its concept). */
#ifndef CT_NARROW_H
#define CT_NARROW_H
#endif
