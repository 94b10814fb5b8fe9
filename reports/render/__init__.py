"""Reports rendered from stored results alone: HTML, Markdown and figures."""
