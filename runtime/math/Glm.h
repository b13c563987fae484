#pragma once

// One place that configures GLM (GLM_FORCE_EXPLICIT_CTOR comes from kiosk_configure_target):
// geodesy and cameras in double, GPU data in float relative to a tile or scene origin.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
