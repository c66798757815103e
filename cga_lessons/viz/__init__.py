"""Drawing: matplotlib 2D/3D figures and the meshcat scene.  Nothing outside viz imports viz."""
