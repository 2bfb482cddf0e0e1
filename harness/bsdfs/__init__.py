"""BSDF conformance: a BSDF's sampling, weights, pdf, energy and reciprocity, at given incident directions."""
