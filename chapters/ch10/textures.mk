CHAPTERS += ch10
ch10_PROGS += ch10_textures
ch10_textures_SRC := chapters/ch10/ch10_textures.c
ch10_textures_MODULES := texture solid noise bumpgen mipmap interp raydiff camera shape cobject frame vec colour image netpbm fileio error
ch10_textures_LIBS := -lm
# what it must not link (make check-links): it shades its pictures
# itself, so no renderer, scene file or image files beyond PPM
ch10_textures_FORBID := render integrator scenefile texpart exrio pngio
