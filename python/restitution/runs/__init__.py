"""Many impacts: sweeps over axes or a cases table (in memory or streamed to a resumable Parquet
dataset), TOML configs, Dask clusters and progress reporting. Uses the scene layer only."""
