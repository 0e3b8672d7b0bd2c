"""Scene: a scenario built in Python with the names of the TOML file (docs/scenario-files.md),
checked by the same reader, so a mistake raises blockdem.ScenarioError (a ValueError) with the
message `blockdem run` prints for the same file."""
import tomllib

from . import _core
from .toml_writer import dumps


class Scene:
    """The tables of a scenario as dicts and lists, in `data`; every method returns the scene so
    that calls chain. Nothing is checked until build() (or to_toml() is read by the engine)."""

    def __init__(self, title=None, file="<python>"):
        self.data = {}
        self.file = file  #: the name errors give as FILE
        if title is not None:
            self.data["title"] = title

    @classmethod
    def from_toml(cls, path):
        """A scene holding a TOML scenario file's tables, to change before build()."""
        with open(path, "rb") as f:
            data = tomllib.load(f)
        scene = cls(file=str(path))
        scene.data = data
        return scene

    @classmethod
    def from_dict(cls, data, file="<python>"):
        scene = cls(file=file)
        scene.data = dict(data)
        return scene

    def _table(self, name, values):
        self.data.setdefault(name, {}).update(values)
        return self

    def _append(self, name, entry):
        self.data.setdefault(name, []).append(entry)
        return self

    # Top-level tables.
    def settings(self, **values):
        """[settings]: gravity, damping, time_step, safety_factor, contact_mode, ..."""
        return self._table("settings", values)

    def output(self, **values):
        """[output]: vtk."""
        return self._table("output", values)

    def voussoir(self, **values):
        """[voussoir]: a voussoir beam (docs/voussoir.md)."""
        return self._table("voussoir", values)

    def rock_mass(self, **values):
        """[rock_mass]: a region cut into blocks by the joint sets (docs/rock-mass.md)."""
        return self._table("rock_mass", values)

    # Arrays of tables.
    def material(self, name, density, **values):
        """[[materials]]: density (kg/m^3)."""
        return self._append("materials", {"name": name, "density": density, **values})

    def joint_law(self, name, normal, shear, **values):
        """[[joint_laws]]: normal = {law, ...}, shear = {law, ..., friction_deg, cohesion, ...}."""
        return self._append("joint_laws", {"name": name, "normal": dict(normal),
                                           "shear": dict(shear), **values})

    def joint(self, groups, law):
        """[[joints]]: the law between blocks of two groups."""
        return self._append("joints", {"groups": list(groups), "law": law})

    def block(self, name, **values):
        """[[blocks]]: any block keys (shape, size, planes, vertices, position, motion, ...)."""
        return self._append("blocks", {"name": name, **values})

    def box(self, name, size, position=(0.0, 0.0, 0.0), **values):
        """A box block of size [lx, ly, lz] (m) centred at position (m)."""
        return self.block(name, shape="box", size=list(size), position=list(position), **values)

    def planes_block(self, name, planes, **values):
        """A block bounded by half-spaces n.x <= d, rows [nx, ny, nz, d]."""
        return self.block(name, shape="planes", planes=[list(p) for p in planes], **values)

    def vertices_block(self, name, vertices, **values):
        """A block as the convex hull of its vertices (m)."""
        return self.block(name, shape="vertices", vertices=[list(v) for v in vertices], **values)

    def joint_set(self, **values):
        """[[joint_sets]] of a rock mass."""
        return self._append("joint_sets", values)

    def excavation(self, name, **values):
        """[[excavations]] of a rock mass."""
        return self._append("excavations", {"name": name, **values})

    def boundary(self, **values):
        """[[boundaries]] of a rock mass."""
        return self._append("boundaries", values)

    def stage(self, name, **values):
        """[[stages]]: kind, gravity, ramp_steps, damping, tolerances, servos, ..."""
        return self._append("stages", {"name": name, **values})

    # Results.
    def to_toml(self):
        """The scene as TOML text (what `blockdem run` would read)."""
        return dumps(self.data)

    def save(self, path):
        """Writes the scene as a TOML file for `blockdem run`."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_toml())

    def build(self):
        """The checked Scenario; raises ScenarioError ('FILE: KEY: REASON')."""
        return _core.Scenario.parse(self.to_toml(), self.file)

    def simulation(self):
        """A Simulation of the built scenario."""
        return _core.Simulation(self.build())
