"""How a user drives FibrilFit inside Blender: scene properties, the sidebar panel, operators
and UI-only scene tools, registered from one list (`registration`). Thin over the same
functions the command line calls."""
