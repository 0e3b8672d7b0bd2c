#!/usr/bin/env python3
"""Writes a three-set rock mass as a blockdem scenario (TOML) for the scale benchmarks.

A cube of rock (side L) cut by three persistent joint sets at 1 m spacing by the [rock_mass]
builder: J1 dip 80 towards 010, J2 dip 75 towards 100, J3 dip 10 towards 230 (three sets at
oblique angles: rhombohedra, and blocks of many shapes at the boundary, not shared cubes).
Sandstone 2500 kg/m^3, linear joints k_n = 5 GPa/m, k_s = 0.5 GPa/m, friction 35 deg, damping 0.7,
automatic time step; no block below 0.0002 m^3 (the cuts that would make
slivers are not made); the base fixed, the sides on rollers; one stage of `steps` steps under
1 g from the blocks as cut (joints exactly closed). L is chosen for about `blocks` blocks before
slivers are avoided (a cube of 1000 m^3 is cut into 1420): --blocks 1000, 10000, 100000 give
L = 8.9, 19.2, 41.3 m and, with the slivers avoided, about 1.0e3, 8.4e3 and 7.6e4 blocks.
With --in-situ the joints start instead with the geostatic stress under 10 m more of rock (the
top carries that traction): the rock mass is at rest from the first step, every joint pressed.

    /usr/bin/python3 bench/make_rockmass.py --blocks 100000 --steps 11 --mode boon2012 > rm.toml
"""
import argparse
import sys


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--blocks", type=int, required=True, help="about this many blocks")
    p.add_argument("--steps", type=int, default=11)
    p.add_argument("--mode", choices=["boon2012", "face_integrated"], default="boon2012")
    p.add_argument("--excavate", type=int, default=0, metavar="STEPS",
                   help="after settling, a stage of STEPS steps that excavates a horseshoe "
                        "tunnel (radius 0.1 L) along y through the cube's middle")
    p.add_argument("--density-scaling", action="store_true",
                   help="density_scaling = true in the stages (quasi-static settling)")
    p.add_argument("--in-situ", action="store_true",
                   help="the joints start with the geostatic stress of 10 m of rock above the "
                        "cube's top (k = 0.5 both ways) and gravity on from the first step: the "
                        "rock mass starts settled, every joint pressed ([in_situ]; the top "
                        "carries the field's traction)")
    p.add_argument("--max-blocks", type=int, default=0,
                   help="[rock_mass] max_blocks (0: the builder's default, 2e6 estimated)")
    a = p.parse_args()
    side = round((a.blocks / 1.42) ** (1.0 / 3.0), 1)
    out = sys.stdout
    out.write(f'title = "three-set rock mass, cube of {side} m, 1 m spacing"\n')
    out.write(f'[settings]\ndamping = 0.7\ncontact_mode = "{a.mode}"\n')
    if a.in_situ:
        out.write("gravity = [0.0, 0.0, -9.81]\n")
    out.write("[output]\nvtk = false\n")
    out.write('[[materials]]\nname = "sandstone"\ndensity = 2500.0\n')
    out.write('[[joint_laws]]\nname = "joint"\nnormal = { law = "linear", stiffness = 5e9 }\n'
              'shear = { law = "linear", stiffness = 5e8, friction_deg = 35 }\n')
    out.write(f'[rock_mass]\nregion = {{ min = [0, 0, 0], max = [{side}, {side}, {side}] }}\n'
              'material = "sandstone"\nlaw = "joint"\n'
              # Slivers at the region's faces are merged into their neighbours (a sliver's
              # half-thickness below the rounding distance is an input error).
              'min_block_volume = 0.0002\n')
    if a.max_blocks > 0:
        out.write(f'max_blocks = {a.max_blocks}\n')
    # The sets pass 0.37 m, 0.61 m and 0.23 m off the region's corner, so no joint runs along a
    # region face.
    for name, dip, direction, origin in (("J1", 80, 10, 0.37), ("J2", 75, 100, 0.61),
                                         ("J3", 10, 230, 0.23)):
        out.write(f'[[joint_sets]]\nname = "{name}"\ndip_deg = {dip}\n'
                  f'dip_direction_deg = {direction}\nspacing = 1.0\n'
                  f'origin = [{origin}, {origin}, {origin}]\nlaw = "joint"\n')
    out.write('[[boundaries]]\nfaces = ["z_min"]\ncondition = "fixed"\n')
    out.write('[[boundaries]]\nfaces = ["x_min", "x_max", "y_min", "y_max"]\n'
              'condition = "roller"\n')
    if a.in_situ:
        out.write(f'[in_situ]\nground_z = {side + 10.0:.1f}\nmaterial = "sandstone"\n'
                  'k_x = 0.5\nk_y = 0.5\n')
        out.write('[[boundaries]]\nfaces = ["z_max"]\ncondition = "stress"\n')
    if a.excavate > 0:
        r = round(0.1 * side, 2)
        out.write(f'[[excavations]]\nname = "tunnel"\nshape = "tunnel"\nprofile = "horseshoe"\n'
                  f'centre = [{side / 2:.2f}, {side / 2:.2f}, {side / 2:.2f}]\nradius = {r}\n'
                  f'wall_height = {r}\ntrend_deg = 0\nplunge_deg = 0\n')
    out.write(f'[[stages]]\nname = "settle"\ngravity = [0.0, 0.0, -9.81]\nkind = "steps"\n'
              f'steps = {a.steps}\n')
    scaling = "density_scaling = true\n" if a.density_scaling else ""
    out.write(scaling)
    if a.excavate > 0:
        out.write(f'[[stages]]\nname = "excavate"\nkind = "steps"\nexcavation = "tunnel"\n'
                  f'steps = {a.excavate}\n{scaling}')


if __name__ == "__main__":
    main()
