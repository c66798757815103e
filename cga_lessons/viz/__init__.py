"""Drawing: matplotlib 2D/3D figures, the notebooks' explorers (widgets) and the meshcat scene.

Layer 5 of the package: imports layers 0-4 only, and nothing below imports it (``tests/test_layers.py`` checks
it).  Its modules are its public face (one per chapter's figures or per explorer), imported by name, e.g.
``from cga_lessons.viz import laser as draw``.
"""

__all__ = [
    "ch2",
    "ch2_3d",
    "ch2_accuracy",
    "ch2_transformations",
    "controls",
    "exploration",
    "explore_conformal_map",
    "explore_entities",
    "explore_motion",
    "explore_nodes",
    "explore_null_cone",
    "explore_products",
    "explore_relocalization",
    "explore_robot",
    "explore_scan",
    "explore_stereo",
    "future_work",
    "future_work_arms",
    "future_work_stereo",
    "future_work_tables",
    "laser",
    "map3d",
    "meshcat_scene",
    "meshcat_server",
    "motions",
    "relocalization",
    "scene3d",
    "scene3d_matplotlib",
    "stereo",
]
