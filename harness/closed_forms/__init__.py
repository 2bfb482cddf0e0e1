"""Scenes whose image is known exactly: a lone plane, a sphere resting on a floor (their geometry and
visibility terms), a furnace; the integrator entries build their closed forms from these."""
