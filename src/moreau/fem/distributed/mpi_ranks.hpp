#pragma once
// The MPI ranks of a distributed run, `mpirun -np N moreau run scene.json`. The engine does not
// link MPI: it learns from the launcher's environment that mpirun started it, and then loads the
// PETSc plugin, which starts MPI and lends the engine its collective operations (Communicator).
// Every rank loads the whole scene and keeps the whole state; the rows of the FEM systems are
// divided among the ranks (mesh_partition.hpp, row_ownership.hpp), rank 0 writes the output.
#include "moreau/fem/petsc/petsc_plugin_api.hpp"

namespace moreau {

/// The number of processes the launcher started: Open MPI's OMPI_COMM_WORLD_SIZE, or PMI_SIZE (MPICH's
/// Hydra, Slurm's PMI); 1 without a launcher.
int launched_ranks();

/// When launched_ranks() > 1: loads the PETSc plugin, which starts MPI. Throws std::runtime_error
/// if the plugin cannot be loaded or MPI's world is not the launcher's.
void start_mpi_if_launched();

/// The ranks of this run, or null on one process (also under `mpirun -np 1`).
const petsc_plugin::Communicator* mpi_world();
/// This process's rank (0 on one process) and the number of ranks (1 on one process).
int mpi_rank();
int mpi_ranks();
/// The largest of `value` over the ranks (`value` itself on one process).
int largest_over_ranks(int value);

}  // namespace moreau
