// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// The saliency detector's building blocks, one header each: MatArena (mat_arena.h), MbdSaliency
// (mbd_saliency.h), RegionExtractor (region_extractor.h) and ExtentGrower (extent_grower.h).
// Included together here for code that uses several of them.
#pragma once

#include "obstacle_tracker/core/extent_grower.h"
#include "obstacle_tracker/core/mat_arena.h"
#include "obstacle_tracker/core/mbd_saliency.h"
#include "obstacle_tracker/core/region_extractor.h"
