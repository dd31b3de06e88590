"""The cell as data: typed scenarios, the plant, frames, object models, the vacuum.

- :mod:`.scenario`: the scenario YAML, loaded typed (misspelled keys refused);
  :mod:`.scenario_sections` the dataclass of each section,
  :mod:`.scenario_checks` the check of each section's values;
  :mod:`.yaml_schema` its strict reader; :mod:`.vacuum` the vacuum key and law.
- :mod:`.plant`: the arm, tool, cell and objects as a ``MultibodyPlant``;
  :mod:`.cup_geometry` the cup's rim spheres and a tool's holders;
  :mod:`.parser` resolves ``package://rt_drake``; :mod:`.frames` the cup
  frame's name and look-up; :mod:`.resources` the shipped files.
- :mod:`.object_model`, :mod:`.object_geometry`, :mod:`.held`: an object's
  model file, its box, and its inertia in the cup frame.
"""
