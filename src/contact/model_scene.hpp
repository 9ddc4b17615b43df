// A contact model's scene side, beside the law and not in it: how a scene names its pair
// coefficients, the example coefficients of `yuxi collide`, and the columns its per-contact
// state gives an analysis. The law's own header (hooke.hpp, linear_spring_dashpot.hpp, ...)
// holds only what runs in the pair loop on any backend (YUXI_HD functions of plain data); each
// model's <model>_scene.hpp specializes ModelScene for it:
//
//   template <class V> static void fields(V& v, Coeffs& c)   the scene keys (scene_fields.hpp)
//   static Coeffs example()                                   in the model units of
//                                                             example_units.hpp
// and optionally
//   static Coeffs with_materials(c, E1, nu1, E2, nu2)         coefficients that also depend on
//                                                             the two materials' elastic
//                                                             constants ([material.<name>])
//   static void lammps_preset(Coeffs& c)                      the defaults of preset = "lammps"
//
// and defines, beside it, `columns(const State&, F&& f)` (state_columns.hpp), which calls
// f(name, value) for each field of the model's state.
#pragma once

namespace yuxi {

template <class Model> struct ModelScene;

} // namespace yuxi
