/* SPDX-License-Identifier: MIT
 * libselftalk umbrella header: everything public. A controller that needs only the network
 * can include selftalk/net.h alone and link libselftalk-core. */
#ifndef SELFTALK_SELFTALK_H
#define SELFTALK_SELFTALK_H

#include "selftalk/base.h"
#include "selftalk/config.h"
#include "selftalk/ga.h"
#include "selftalk/genome.h"
#include "selftalk/io.h"
#include "selftalk/net.h"
#include "selftalk/rng.h"

#endif
