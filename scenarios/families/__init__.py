"""The mechanism families, one module each; each declares itself as a `Family` (scenarios/family.py)."""
