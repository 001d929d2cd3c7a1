"""Syntax to description: the XML frontend and the substitution tokenizer."""
