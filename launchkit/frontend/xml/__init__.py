"""The XML frontend: lxml elements with file:line:col, parsed into the description."""
