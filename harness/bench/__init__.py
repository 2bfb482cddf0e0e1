"""Speed against error: sample-count ladders for each engine and their reports."""
