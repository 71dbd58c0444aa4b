// glTF alpha coverage, shared by the G-buffer and the shadow passes: the factor times the
// vertex alpha times the texture's alpha at full resolution (textureLod 0), the texels the
// ground truth's CPU test (Scene::coverage) reads. Mipmapped alpha would thin foliage out with
// distance and differ between the camera's and the light's views.
#ifndef PENUMBRA_ALPHA_TEST_GLSL
#define PENUMBRA_ALPHA_TEST_GLSL

// `alphaTest`, `hasTexture`: the material's flags, or the G-buffer's specialization constants
// (lavapipe samples a texture under a false branch all the same).
bool coverageHole(MaterialPush m, sampler2D baseColorTexture, vec2 uv, float vertexAlpha,
                  bool alphaTest, bool hasTexture) {
    if (!alphaTest) return false;
    float alpha = m.baseColor.a * vertexAlpha;
    if (hasTexture) alpha *= textureLod(baseColorTexture, uv, 0.0).a;
    return alpha < m.alphaCutoff;
}

#endif
