CHAPTERS += ch06
ch06_PROGS += ch06_display
ch06_display_SRC := chapters/ch06/ch06_display.c
ch06_display_MODULES := tonemap image netpbm fileio colour error
ch06_display_LIBS := -lm
