/* SPDX-License-Identifier: MIT
 * libselftalk umbrella header: everything public. A controller that needs only the network
 * can include selftalk/net.h alone and link libselftalk-core. */
#ifndef SELFTALK_SELFTALK_H
#define SELFTALK_SELFTALK_H

#include "selftalk/assemble.h"
#include "selftalk/base.h"
#include "selftalk/config.h"
#include "selftalk/csv.h"
#include "selftalk/ga.h"
#include "selftalk/genome.h"
#include "selftalk/io.h"
#include "selftalk/net.h"
#include "selftalk/prediction.h"
#include "selftalk/rng.h"
#include "selftalk/stats.h"
#include "selftalk/study.h"
/* the simulator side (links ODE, urdfdom, assimp): robot, world, sensors, stages */
#include "selftalk/caretaker.h"
#include "selftalk/episode.h"
#include "selftalk/evolve.h"
#include "selftalk/fitnesscsv.h"
#include "selftalk/fitness.h"
#include "selftalk/ik.h"
#include "selftalk/integrated.h"
#include "selftalk/model.h"
#include "selftalk/postcsv.h"
#include "selftalk/posteval.h"
#include "selftalk/poststats.h"
#include "selftalk/postures.h"
#include "selftalk/robot.h"
#include "selftalk/scene.h"
#include "selftalk/scripted.h"
#include "selftalk/sensors.h"
#include "selftalk/trial.h"
#include "selftalk/trialkind.h"
#include "selftalk/world.h"

#endif
