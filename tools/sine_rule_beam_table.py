#!/usr/bin/env python3
"""Writes a sonarsim beam table (assets/devices/beam_tables/*.csv) for a sonar whose beams are evenly spaced in
sin(bearing): centre_i = asin(sin(H) * (1 - 2 i / (N - 1))), i = 0 .. N - 1, beam 0 at +H (port). Edges are the
midpoints between neighbouring centres, the outer ones half a spacing beyond the last centre. The rule is the
one Tritech Gemini and Blueprint Oculus heads report (see the header each table gets); nothing is copied.

Usage: tools/sine_rule_beam_table.py NAME HALF_APERTURE_DEG BEAMS "TITLE" "SOURCE" "CONVENTION" > FILE
"""
import math
import sys


def main(argv):
    if len(argv) != 7:
        sys.stderr.write(__doc__)
        return 2
    _, name, half_deg, beams, title, source, convention = argv
    h, n = math.radians(float(half_deg)), int(beams)
    centres = [math.degrees(math.asin(math.sin(h) * (1 - 2 * i / (n - 1)))) for i in range(n)]
    edges = [centres[0] + (centres[0] - centres[1]) / 2]
    edges += [(centres[i] + centres[i + 1]) / 2 for i in range(n - 1)]
    edges += [centres[-1] - (centres[-2] - centres[-1]) / 2]
    out = sys.stdout
    out.write(f"# sonarsim beam table: {title}\n")
    out.write(f"# source: {source}\n")
    out.write("# licence: numbers computed here from the rule by tools/sine_rule_beam_table.py (no table copied)\n")
    out.write(f"# convention: {convention}\n")
    out.write("# columns: beam (sonarsim, 0 = port-most), device_beam (the device's own number), centre_deg, "
              "port_edge_deg, starboard_edge_deg [deg, positive = port], gain (relative response, 1 = none)\n")
    out.write("beam,device_beam,centre_deg,port_edge_deg,starboard_edge_deg,gain\n")
    for i in range(n):
        out.write(f"{i},{i},{centres[i]:.6f},{edges[i]:.6f},{edges[i + 1]:.6f},1\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
