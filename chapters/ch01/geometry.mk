CHAPTERS += ch01
ch01_PROGS += ch01_geometry
ch01_geometry_SRC := chapters/ch01/ch01_geometry.c
ch01_geometry_MODULES := vec frame ray bbox cobject error shape quadric sphere plane disk parallelogram triangle box cylinder cone xform camera
ch01_geometry_LIBS := -lm
