// sss-render's float simulators (render.precision = "float"): the whitelist's float instantiations, and the
// seabed's synthesis, float in both scalars (scene_file/build.hpp, make_seabed).
#include "render_scene.hpp"

template int sss::scene_file::render_scene<float>(const sss::scene_file::description&, const sss::scene_file::render_request&);
template sss::seabed::composite_seabed<float> sss::scene_file::synthesise_seabed<float>(const sss::scene_file::description&);
