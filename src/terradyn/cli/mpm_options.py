"""The options shared by the ``terradyn mpm`` commands (one definition each)."""

from __future__ import annotations

import typer


class MPMOptions:
    cell_size = typer.Option(
        None, "--cell-size", help="Grid cell size [m] (default: diameter / 20, wheels / 32)."
    )
    ppc = typer.Option(2, "--particles-per-cell", help="Particles per cell along each axis.")
    volumetric = typer.Option(
        "point",
        "--volumetric",
        help="Velocity divergence of the volume and stress update: point (each point its own, the classical "
        "update) or patch (averaged over the points of a cell, against volumetric locking; docs/mpm.md).",
    )
    flip = typer.Option(
        0.0,
        "--flip",
        help="FLIP fraction of the grains' velocity update, 0-1 (0: APIC alone). APIC's numerical viscosity "
        "raises forces with speed / cfl at the cell scale; 0.99 removes most of it (docs/mpm.md, 'What the "
        "rate error is').",
    )
    packing = typer.Option("consolidated", "--packing", help="consolidated or unconsolidated bed.")
    walls = typer.Option(None, "--walls", help="Wall condition: free-slip, no-slip or frictional.")
    contact = typer.Option(
        "two-field",
        "--contact",
        help="Body-grain grid contact: two-field (default), two-field-gap (contact once the grains reach "
        "the body, docs/mpm.md 'Contact at a distance') or the legacy cover.",
    )
    checkpoint = typer.Option(
        None, "--checkpoint", help="Checkpoint file (.npz), written atomically, on Ctrl-C and at the end."
    )
    checkpoint_interval = typer.Option(
        60.0, "--checkpoint-interval", help="Wall-clock seconds [s] between checkpoints."
    )
    resume = typer.Option(False, "--resume", help="Continue the run saved in --checkpoint (it must exist).")
    snapshots = typer.Option(
        None, "--snapshots", help="Folder for particle snapshots (NetCDF, fields extra)."
    )
    series = typer.Option(None, "--series", help="Time series file (.csv).")
    fields = typer.Option(
        None, "--fields", help="Particle speed and pressure at the end of the run (.png/.pdf/.svg/.jpg)."
    )
    frames = typer.Option(40, "--frames", help="Frames in the --animate animation (2-500).")
    record_interval = typer.Option(
        None,
        "--record-interval",
        help="Simulated time [s] per time-series row (default: a quarter cell of travel).",
    )
    snapshot_interval = typer.Option(
        None,
        "--snapshot-interval",
        help="Simulated time [s] between --snapshots files (default: 4 cells of travel).",
    )
    plot = typer.Option(None, "--plot", help="Force history plot (.png/.pdf/.svg/.jpg).")
    dilatancy = typer.Option(
        0.0,
        "--dilatancy",
        help="Dilatancy coefficient K [-] of tan(psi) = K (phi - phi_c): dense beds dilate, loose ones "
        "compact and stay as loose as prepared; 0 = off (isochoric flow).",
    )
    surface_friction = typer.Option(
        None,
        "--surface-friction",
        help="Body-grain Coulomb friction [-] (0-2; default: the medium's, 0.4 in the shipped ones). "
        "It limits a wheel's thrust: calibrate it with the bed before comparing pulls (docs/mpm.md).",
    )
