CHAPTERS += ch07
ch07_PROGS += ch07_grids
ch07_grids_SRC := chapters/ch07/ch07_grids.c
ch07_grids_MODULES := accel grid grid_build primset mesh meshgen triangle shape frame vec bbox cobject ray rng error camera image netpbm fileio
ch07_grids_LIBS := -lm
# what it must not link (make check-links): its scenes are meshes alone,
# so no parallelogram, transform, batched brute force, renderer, photon
# map or texture
ch07_grids_FORBID := volphoton parallelogram xform batch render integrator tracer photon irrpart irrcache gradients texture texpart noise_ solid_ mipmap bumpgen interp_
