// The "W" shape of the spanwise profile (seed paper section 4.4, Fig. 15(b)): at mid-stroke the
// dorsal and ventral edges lead and the middle of the fin lags. Per half of the spanwise line
// (1 = dorsal/upper, 2 = ventral/lower): d is the lateral distance from the convex region (the
// edge tip) to the concave region (the node of that half lagging furthest behind the tip), and
// alpha the angle to the vertical of the line joining them. The paper's values: reconstruction
// alpha1 41 deg, alpha2 32 deg, d1 0.086c, d2 0.165c; its FSI 40 deg, 19 deg, 0.060c, 0.126c.
// "Behind" is the side opposite to where the two tips' mean sits relative to mid-span, so the
// measure does not depend on the stroke's direction. A half with no lag gives d = 0, alpha = 0.
#pragma once

#include <vector>

namespace finverse::report {

struct WShape {
  double alpha1_deg = 0, alpha2_deg = 0;  // upper, lower half
  double d1 = 0, d2 = 0;                  // in chords
};

// z: spanwise coordinate of the line's nodes, ascending [m]; y: their lateral position [m];
// chord [m]. Throws finverse::Error for fewer than 3 nodes, unsorted z or mismatched sizes.
WShape w_shape(const std::vector<double>& z, const std::vector<double>& y, double chord);

}  // namespace finverse::report
