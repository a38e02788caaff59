#pragma once
//! The element-wise N_Vector operations CVODE runs on the state vector, compiled with the
//! project (optimised).
//!
//! Debian 12's SUNDIALS 6.4.1 is built without optimisation (its N_VLinearSum_Serial
//! keeps its loop counter on the stack: `objdump -d libsundials_cvode.so.6.4.1`), so the
//! vector kernels of every BDF step, Newton iteration and error test ran several times
//! slower than they need to (tests/bench/README.md, Performance).
//! install_serial_vector_ops() points a serial vector's operation table at the functions
//! below; CVODE clones its work vectors from the state vector, operations included. Each
//! function does exactly the arithmetic of the library's (the same special cases where
//! they round differently: a (x + y) for N_VLinearSum with a == b, a (x - y) with a ==
//! -b), so a run gives the same bits; `SerialVectorOps.*` compares every one with the
//! library's, bit for bit.
#include <nvector/nvector_serial.h>

namespace panoptic {

void install_serial_vector_ops(N_Vector v);

}  // namespace panoptic
