"""Cube configs: the TOML file of `gradem specimen`, `compress` and `tension`, with typed overrides.

An override is the key written into the config's TOML document, which the config reader then
reads again: the names, units, defaults, ranges and messages are the file's
(experiments/README.md "Config keys"). A refused value raises gradem.InputError (a ValueError)
naming the key, the value and the allowed values, and leaves the config as it was.

    cfg = gradem.CubeConfig.load("experiments/configs/calibration_cube.toml")
    cfg.material.tensile_strength_mpa = 12        # [material] keys: the material table's rows
    cfg.genesis.edge_mm = 2.0                     # any other key of the file
    cfg["test.stop_fraction"] = 0.8               # the same, by name
    del cfg.material.cohesion_mpa                 # back to the default
    cfg.set({"material.model": "soft_bond", "material.softening_factor": 0.2})  # together
    sweep = [cfg.copy({"material.tensile_strength_mpa": s}) for s in (8, 10, 12)]
    cfg.save("my_cube.toml")                      # `gradem compress my_cube.toml` runs the same test
"""

import os

from . import _gradem

# The tables of an explicit-paste config, which a parallel-bond config does not list.
_PASTE_TABLES = ("mix", "paste")


def material_table():
    """Every [material] key: its unit, type, allowed range, the bond models it belongs to."""
    return _gradem.material_table()


class _Section:
    """One [table] of a config: its keys as attributes (read and set)."""

    __slots__ = ("_config", "_table")

    def __init__(self, config, table):
        object.__setattr__(self, "_config", config)
        object.__setattr__(self, "_table", table)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return self._config[f"{self._table}.{name}"]

    def __setattr__(self, name, value):
        self._config.set({f"{self._table}.{name}": value})

    def __delattr__(self, name):
        self._config.set({f"{self._table}.{name}": None})

    def __getitem__(self, name):
        return self._config[f"{self._table}.{name}"]

    def __setitem__(self, name, value):
        self._config.set({f"{self._table}.{name}": value})

    def keys(self):
        if self._table == "material":
            return list(self._config._impl.material_keys)
        prefix = self._table + "."
        return [k[len(prefix):] for k in self._config._impl.keys() if k.startswith(prefix)]

    def __dir__(self):
        return self.keys()

    def to_dict(self):
        return {k: self[k] for k in self.keys()}

    def __repr__(self):
        rows = "".join(f"\n  {k} = {v!r}" for k, v in self.to_dict().items())
        return f"[{self._table}]{rows}"


class CubeConfig:
    """A cube config (experiments/README.md): load(), typed overrides, save()."""

    __slots__ = ("_impl",)

    def __init__(self, impl):
        object.__setattr__(self, "_impl", impl)

    @classmethod
    def load(cls, path):
        """Reads and checks a cube config TOML file (gradem.InputError naming file, line and key)."""
        return cls(_gradem.Config.load(os.fspath(path)))

    @property
    def file(self):
        """The TOML file it was loaded from (paths in it are relative to its folder)."""
        return self._impl.file

    @property
    def bond_model(self):
        return self._impl.bond_model

    @property
    def overrides(self):
        """The keys set since load(), as TOML values ("(default)": removed)."""
        return dict(self._impl.overrides)

    def _tables(self):
        tables = {k.split(".", 1)[0] for k in self._impl.keys()}
        return sorted(tables | {"material", "tension"})

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._tables() or name in _PASTE_TABLES:
            return _Section(self, name)
        raise AttributeError(f"CubeConfig has no attribute or table '{name}' (tables: {', '.join(self._tables())})")

    def __setattr__(self, name, value):
        raise AttributeError(f"set a key of a table, e.g. cfg.material.tensile_strength_mpa = 12 (not cfg.{name})")

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._tables()))

    def __getitem__(self, key):
        """The value of 'table.key' in config units (its default when the file does not give it)."""
        return self._impl.get(key)

    def __setitem__(self, key, value):
        self.set({key: value})

    def __delitem__(self, key):
        self.set({key: None})

    def set(self, overrides):
        """Sets several keys at once ({'table.key': value, ...}; None: the default): all or none."""
        self._impl.set(dict(overrides))
        return self

    def copy(self, overrides=None):
        """A copy, with `overrides` ({'table.key': value}) applied to it."""
        c = CubeConfig(self._impl.copy())
        if overrides:
            c.set(overrides)
        return c

    def keys(self):
        """Every key the reader knows, 'table.key' -> value (config units)."""
        return {k: row["value"] for k, row in self._impl.keys().items()}

    def describe(self):
        """Every key: value, the line that gives it (0: the default or an override) and whether it is a path."""
        return self._impl.keys()

    def document(self):
        """The TOML document as it stands (the file with the overrides)."""
        return self._impl.document()

    def save(self, path):
        """Writes the config as TOML (paths absolute, comments dropped), atomically."""
        self._impl.save(os.fspath(path))

    def __repr__(self):
        extra = f", overrides={self.overrides}" if self.overrides else ""
        return f"CubeConfig({self.file!r}{extra})"


def as_impl(config):
    """The extension's config of a CubeConfig or a path."""
    if isinstance(config, CubeConfig):
        return config._impl
    if isinstance(config, (str, os.PathLike)):
        return _gradem.Config.load(os.fspath(config))
    raise TypeError(f"expected a gradem.CubeConfig or the path of a cube config, got {type(config).__name__}")
