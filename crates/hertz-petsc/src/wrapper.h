/* Everything hertz-petsc calls lives behind petscksp.h (petscmat.h, petscvec.h, petscsys.h, mpi.h). */
#include <petscksp.h>
