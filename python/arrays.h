#pragma once
// NumPy views of results Penumbra already holds: no copy. Each array keeps the C++ result alive
// through a capsule, so the pixels live as long as any array (or the result object) does.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

namespace penumbra::python {

namespace py = pybind11;

// An array over `data` (C order, `shape`), owned by `owner`; writes go to the result itself, so
// metrics() sees whatever the caller changed.
template <class T, class Owner>
py::array_t<T> viewOf(std::vector<T>& data, std::vector<py::ssize_t> shape,
                      const std::shared_ptr<Owner>& owner) {
    auto* keep = new std::shared_ptr<Owner>(owner);
    py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Owner>*>(p); });
    return py::array_t<T>(std::move(shape), data.data(), base);
}

// One (height, width) array per image of `images` (a light's visibility, its occluder distance).
template <class Owner>
py::list viewsOf(std::vector<std::vector<float>>& images, uint32_t width, uint32_t height,
                 const std::shared_ptr<Owner>& owner) {
    py::list out;
    for (std::vector<float>& image : images)
        out.append(viewOf(image, {py::ssize_t(height), py::ssize_t(width)}, owner));
    return out;
}

// One (height, width, 3) array per image of `images` (a light's light per channel, linear RGB).
template <class Owner>
py::list rgbViewsOf(std::vector<std::vector<float>>& images, uint32_t width, uint32_t height,
                    const std::shared_ptr<Owner>& owner) {
    py::list out;
    for (std::vector<float>& image : images)
        out.append(viewOf(image, {py::ssize_t(height), py::ssize_t(width), py::ssize_t(3)}, owner));
    return out;
}

} // namespace penumbra::python
