// sss-render's double simulators (render.precision = "double"): the whitelist's double instantiations.
#include "render_scene.hpp"

template int sss::scene_file::render_scene<double>(const sss::scene_file::description&, const sss::scene_file::render_request&);
