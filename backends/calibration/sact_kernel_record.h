#pragma once
#include "robocore/collision/sact_kernel_record.h"  // moved to robocore (the RoboCore API's CheckCollisions)
