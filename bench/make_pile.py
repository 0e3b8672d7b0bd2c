#!/usr/bin/env python3
"""Writes a 3D running-bond brick pile as a blockdem scenario (TOML) for the scale benchmarks.

Layout (the pile of the performance audit): 46 mm gypsum cubes (1207 kg/m^3) on a fixed base
plate; even layers n x n cubes, odd layers (n-1) x (n-1) shifted by half a cube in x and y, each
resting on four below; layers pre-closed by 50 nm; side faces exactly touching. Linear joints
k_n = 10 GPa/m, k_s = 1 GPa/m, friction 40 deg, damping 0.7, automatic time step, one stage of
`steps` steps under 1 g, no VTK output.

    /usr/bin/python3 bench/make_pile.py --n 100 --layers 10 --steps 11 --mode boon2012 > pile.toml
"""
import argparse
import sys


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, required=True, help="cubes per side of an even layer")
    p.add_argument("--layers", type=int, default=10)
    p.add_argument("--steps", type=int, default=11)
    p.add_argument("--mode", choices=["boon2012", "face_integrated"], default="boon2012")
    a = p.parse_args()
    s, pre = 0.046, 5e-8
    out = sys.stdout
    out.write(f'title = "running-bond brick pile n={a.n} layers={a.layers}"\n')
    out.write(f'[settings]\ndamping = 0.7\ncontact_mode = "{a.mode}"\n')
    out.write("[output]\nvtk = false\n")
    out.write('[[materials]]\nname = "gypsum"\ndensity = 1207.0\n')
    out.write('[[joint_laws]]\nname = "joint"\nnormal = { law = "linear", stiffness = 10e9 }\n'
              'shear = { law = "linear", stiffness = 1e9, friction_deg = 40 }\n')
    w = (a.n + 2) * s
    out.write(f'[[blocks]]\nname = "base"\nmaterial = "gypsum"\nsize = [{w}, {w}, {s}]\n'
              f'position = [{0.5 * a.n * s}, {0.5 * a.n * s}, {-0.5 * s}]\nmotion = "fixed"\n')
    k = 0
    for layer in range(a.layers):
        m = a.n if layer % 2 == 0 else a.n - 1
        shift = 0.0 if layer % 2 == 0 else 0.5 * s
        z = (layer + 0.5) * s - (layer + 1) * pre
        for i in range(m):
            for j in range(m):
                out.write(f'[[blocks]]\nname = "c{k}"\nmaterial = "gypsum"\n'
                          f'size = [{s}, {s}, {s}]\n'
                          f'position = [{shift + (i + 0.5) * s!r}, {shift + (j + 0.5) * s!r}, {z!r}]\n')
                k += 1
    out.write(f'[[stages]]\nname = "settle"\ngravity = [0.0, 0.0, -9.81]\nkind = "steps"\n'
              f'steps = {a.steps}\n')


if __name__ == "__main__":
    main()
