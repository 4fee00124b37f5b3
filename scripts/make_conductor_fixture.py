#!/usr/bin/env python3
"""Writes tests/data/conductor_spectra.txt, the spectra the conductor-table test converts on its own.

Usage: python3 scripts/make_conductor_fixture.py MITSUBA_DATA_DIR > tests/data/conductor_spectra.txt

Each of mitsuba-data's ior/NAME.{eta,k}.spd tables (see scripts/make_conductors.py for their
sources) restricted to 360-830 nm: the table's own points there, and its values at every 5 nm
in that span inside the table's range (so that the span's ends interpolate as the full table does). One line per table:
NAME eta|k  wavelength:value ...
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_conductors as mc  # noqa: E402


def main():
    ior, names = mc.tables(sys.argv, __doc__)
    print("# Resampled by scripts/make_conductor_fixture.py from mitsuba-data's ior/ tables")
    print("# (luxpop.com, after Palik's Handbook of Optical Constants of Solids). nm:value")
    for name in names:
        for part in ("eta", "k"):
            pairs = mc.read_spd(os.path.join(ior, "%s.%s.spd" % (name, part)))
            lo, hi = pairs[0][0], pairs[-1][0]
            at = sorted({l for l, _ in pairs if 360.0 <= l <= 830.0} |
                        {360.0 + 5.0 * i for i in range(95) if lo <= 360.0 + 5.0 * i <= hi})
            print(name, part, " ".join("%.6g:%.6g" % (l, mc.value_at(pairs, l)) for l in at))


if __name__ == "__main__":
    main()
