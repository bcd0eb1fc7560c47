// `mpirun -n N relume ...`: when the process was started by mpirun (OpenMPI's or a PMI
// launcher's environment), it joins MPI_COMM_WORLD and installs its ranks for the library
// (core/ranks.hpp), over which a streamed compression splits its pixel rows. Built only with MPI
// (CMake option RELUME_MPI, on when MPI is found); otherwise relume always runs as one process.
#pragma once

namespace relume {

class MpiRun {
 public:
  // Joins the job when started by mpirun; else does nothing (one process).
  MpiRun(int* argc, char*** argv);
  ~MpiRun();  // MPI_Finalize
  MpiRun(const MpiRun&) = delete;
  MpiRun& operator=(const MpiRun&) = delete;

  bool several() const;  // more than one rank
  int rank() const;
  int size() const;
  // Ends every rank with `code` (MPI_Abort): after one rank fails, the others would otherwise wait
  // for it forever in their next exchange.
  [[noreturn]] void abort_all(int code);

 private:
  bool joined_ = false;
};

}  // namespace relume
