/* ct_assemble.h -- part of contact.h (to be filled by its concept). */
#ifndef CT_ASSEMBLE_H
#define CT_ASSEMBLE_H
#endif
