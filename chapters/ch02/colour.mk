CHAPTERS += ch02
ch02_PROGS += ch02_colour
ch02_colour_SRC := chapters/ch02/ch02_colour.c
ch02_colour_MODULES := colour spectrum error
ch02_colour_LIBS := -lm
