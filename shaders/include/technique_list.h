// The technique list, read by C++ and by GLSL: one line per technique, the only place that
// enumerates them. Every reader defines PENUMBRA_TECHNIQUE(id, Name, module, shader) before
// including this file and gets it undefined after:
//   id      the value of penumbra::Technique::Name (include/penumbra/settings.h) and of the
//           visibility pass's TECHNIQUE specialization constant
//   Name    the enum value, and the suffix of the technique's GLSL entry point
//           `vec4 evaluate<Name>(TechniqueInput at)` (shaders/include/techniques.glsl)
//   module  its module, `const TechniqueModule& <module>Module()` (src/shadows/technique.h),
//           which holds everything else: name, parameters, maps, passes, capabilities, packing
//           and CPU reference
//   shader  the GLSL include (shaders/include/<shader>.glsl) that defines evaluate<Name>; the
//           build includes each named file once into techniques.glsl (cmake/Shaders.cmake
//           writes technique_shaders.glsl), so several techniques may share one
// The order is `penumbra techniques`' order. Adding a technique: docs/architecture.md.
// (No include guard: each reader expands it its own way.)
//
// Two roles, named here so that no shared file names a technique (include/penumbra/settings.h):
//   PENUMBRA_DEFAULT_TECHNIQUE   what every command, the Python module and a benchmark run use
//                                when none is named: the plain depth test, the reference point
//                                every other technique is measured against
//   PENUMBRA_COMPARED_TECHNIQUE  the viewer's technique B in its A/B split when none is named
#ifndef PENUMBRA_DEFAULT_TECHNIQUE
#define PENUMBRA_DEFAULT_TECHNIQUE Hard
#define PENUMBRA_COMPARED_TECHNIQUE Pcss
#endif
PENUMBRA_TECHNIQUE(0, Hard, hard, shadow_hard)
PENUMBRA_TECHNIQUE(1, Pcf, pcf, shadow_pcf)
PENUMBRA_TECHNIQUE(2, Pcss, pcss, shadow_pcss)
PENUMBRA_TECHNIQUE(3, SecondDepth, secondDepth, shadow_second_depth)
PENUMBRA_TECHNIQUE(4, Vsm, vsm, shadow_moments)
PENUMBRA_TECHNIQUE(5, Esm, esm, shadow_moments)
PENUMBRA_TECHNIQUE(6, Evsm, evsm, shadow_moments)
PENUMBRA_TECHNIQUE(7, Savsm, savsm, shadow_sat)
PENUMBRA_TECHNIQUE(8, Msm, msm, shadow_moments)
PENUMBRA_TECHNIQUE(9, Vssm, vssm, shadow_sat)
PENUMBRA_TECHNIQUE(10, MsmSoft, msmSoft, shadow_sat)
PENUMBRA_TECHNIQUE(11, Sdf, sdf, shadow_sdf)
PENUMBRA_TECHNIQUE(12, Smrt, smrt, shadow_smrt)
#undef PENUMBRA_TECHNIQUE
