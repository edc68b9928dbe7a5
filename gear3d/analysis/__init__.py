"""Independent checks: brute-force cutting simulation, pair rolling, comparisons."""
