"""Reports: terminal tables, HTML pages and plots. Only this package formats; only the CLI prints."""
