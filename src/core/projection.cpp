#include "core/projection.h"

#include <cmath>

namespace penumbra {

glm::mat4 lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
    const glm::vec3 back = glm::normalize(eye - target); // view +Z
    const glm::vec3 right = glm::normalize(glm::cross(up, back));
    const glm::vec3 trueUp = glm::cross(back, right);
    glm::mat4 m(1.0f);
    for (int i = 0; i < 3; ++i) {
        m[i][0] = right[i];
        m[i][1] = trueUp[i];
        m[i][2] = back[i];
    }
    m[3] = glm::vec4(-glm::dot(right, eye), -glm::dot(trueUp, eye), -glm::dot(back, eye), 1.0f);
    return m;
}

// x' = (2x - (r + l)) / (r - l); y' likewise; depth g(-z) = a(-z) + b with g(n) = 0, g(f) = 1,
// so a = 1/(f - n), b = -n/(f - n). The seeds' last row (row-vector form) is therefore
// [0, 0, n/(n - f), 1]: their printed 2/h in it is a typo.
glm::mat4 orthographic(float l, float r, float b, float t, float n, float f) {
    glm::mat4 m(0.0f);
    m[0][0] = 2.0f / (r - l);
    m[1][1] = 2.0f / (t - b);
    m[2][2] = -1.0f / (f - n);
    m[3][0] = -(r + l) / (r - l);
    m[3][1] = -(t + b) / (t - b);
    m[3][2] = -n / (f - n);
    m[3][3] = 1.0f;
    return m;
}

// w_clip = -z; depth = (A z + B) / (-z) must be 0 at -z = n and 1 at -z = f:
// A = -f/(f - n), B = -f n/(f - n).
glm::mat4 perspectiveLight(float yfov, float aspect, float n, float f) {
    const float cot = 1.0f / std::tan(0.5f * yfov);
    glm::mat4 m(0.0f);
    m[0][0] = cot / aspect;
    m[1][1] = cot;
    m[2][2] = -f / (f - n);
    m[2][3] = -1.0f;
    m[3][2] = -f * n / (f - n);
    return m;
}

// Reverse-Z: depth = (A z + B)/(-z) with 1 at -z = n and 0 at -z = f: A = n/(f - n),
// B = f n/(f - n). y is negated so that +Y (up) lands on the framebuffer's first rows.
glm::mat4 perspectiveCameraReverseZ(float yfov, float aspect, float n, float f) {
    const float cot = 1.0f / std::tan(0.5f * yfov);
    glm::mat4 m(0.0f);
    m[0][0] = cot / aspect;
    m[1][1] = -cot;
    m[2][2] = n / (f - n);
    m[2][3] = -1.0f;
    m[3][2] = f * n / (f - n);
    return m;
}

// depth(t) = (f - t) / (f - n) for distance t = -z: 1 at n, 0 at f.
glm::mat4 orthographicCameraReverseZ(float ymag, float aspect, float n, float f) {
    glm::mat4 m(0.0f);
    m[0][0] = 1.0f / (ymag * aspect);
    m[1][1] = -1.0f / ymag;
    m[2][2] = 1.0f / (f - n);
    m[3][2] = f / (f - n);
    m[3][3] = 1.0f;
    return m;
}

glm::mat4 textureMatrix() {
    glm::mat4 m(1.0f);
    m[0][0] = 0.5f;
    m[1][1] = 0.5f;
    m[3][0] = 0.5f;
    m[3][1] = 0.5f;
    return m;
}

glm::mat4 cameraProjection(const Camera& camera, float aspect) {
    return camera.orthographic
               ? orthographicCameraReverseZ(camera.ymag, aspect, camera.znear, camera.zfar)
               : perspectiveCameraReverseZ(camera.yfov, aspect, camera.znear, camera.zfar);
}

glm::mat4 cameraViewProj(const Camera& camera, float aspect) {
    return cameraProjection(camera, aspect) * lookAt(camera.position, camera.target, camera.up);
}

} // namespace penumbra
