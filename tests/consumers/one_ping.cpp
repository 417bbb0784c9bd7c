#include <sss/sss.hpp>
int main() {
    sss::simulator<> sim;                       // default policies, double
    sss::scene::flat_seabed<double> seabed;     // z = 0
    const auto lines = sim.ping(seabed, 0);     // one ping: lines.port, lines.starboard (std::vector<double>)
    double e = 0; for (double v : lines.starboard) e += v;
    return (lines.port.size() == lines.starboard.size() && e > 0) ? 0 : 1;
}
