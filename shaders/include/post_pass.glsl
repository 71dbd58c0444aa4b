// What every shadow-map post pass that reads its view binds: the view records and the push block
// (PostPassPush.size.z: the view's index). A pass that reads its technique's parameters includes
// the technique's parameter block (TECH_PARAMS) too.
// Inputs and outputs are the pass's own (POST_INPUT_BINDING + i, POST_OUTPUT_BINDING + i).
#ifndef PENUMBRA_POST_PASS_GLSL
#define PENUMBRA_POST_PASS_GLSL
#include "light_geometry.h"
#include "bindings.h"
#include "pass_types.h"
layout(set = 0, binding = POST_VIEWS_BINDING, std140) uniform Views {
    ShadowViewData views[MAX_UNIFORM_VIEWS];
};
layout(push_constant) uniform Push { PostPassPush push; };
#endif
