// The kernel body built for the instruction set named in CMakeLists.txt's flags for this file.
#define PCB_KERNEL_VARIANT avx512
#include "BilateralKernelBody.h"
#include "EdgeAwareKernelBody.h"
