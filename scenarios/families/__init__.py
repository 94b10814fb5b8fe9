"""Mechanism families, one module each."""
