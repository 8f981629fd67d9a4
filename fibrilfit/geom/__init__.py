"""Plain geometry on numpy arrays, no bpy: core outlines and polygons (`polygons`), rigid-body
superposition and screw axes (`rigid`)."""
