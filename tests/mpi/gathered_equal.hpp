// For the MPI tests: a field on the ranks' blocks, gathered onto rank 0, against the serial
// field on the whole grid, bit for bit; the first three differing cells are reported.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "cfd/parallel/distributed_grid.hpp"

inline void expect_gathered_equal(const finverse::cfd::DistributedGrid& g, const finverse::cfd::Field& local,
                                  const finverse::cfd::Field& serial, const std::string& what) {
  finverse::cfd::Field gathered(serial.nx(), serial.ny(), serial.nz(), serial.dim(), 0);
  g.gather(local, gathered);
  if (g.rank() != 0) return;
  int wrong = 0;
  for (int k = 0; k < serial.nz(); ++k)
    for (int j = 0; j < serial.ny(); ++j)
      for (int i = 0; i < serial.nx(); ++i)
        if (gathered(i, j, k) != serial(i, j, k) && ++wrong <= 3)
          ADD_FAILURE() << what << " at (" << i << "," << j << "," << k << "): " << gathered(i, j, k) << " on " << g.size()
                        << " ranks, " << serial(i, j, k) << " serial";
  EXPECT_EQ(wrong, 0) << what;
}
