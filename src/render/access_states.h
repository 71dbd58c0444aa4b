#pragma once
// What each Access means to the device (render/resource_pool.h): the stages, accesses and image
// layout a barrier waits on or moves to, and whether a use writes or reads what it finds.
#include "render/resource_pool.h"
#include "vk/sync.h"

namespace penumbra::render {

vk::ImageState imageState(Access access);   // fatal for a buffer's access
vk::BufferState bufferState(Access access); // fatal for an image's access

} // namespace penumbra::render
