# SPDX-License-Identifier: MIT
"""One key of a run's config.ini (./apps/evolve writes every key under its [section]), for the
tools that read a run directory: the one reader of it they share."""
import os


def value(run_dir, section, key, default, conv):
    """section.key of RUN_DIR/config.ini converted by conv (int, float), default when the
    directory has no config.ini or the file no such key; a value conv refuses raises
    ValueError naming FILE:LINE, the key and what was expected"""
    path = os.path.join(run_dir, "config.ini")
    current = None
    try:
        with open(path) as f:
            for n, line in enumerate(f, start=1):
                line = line.split("#")[0].split(";")[0].strip()
                if line.startswith("["):
                    current = line.strip("[]").strip()
                elif current == section and "=" in line and line.split("=", 1)[0].strip() == key:
                    text = line.split("=", 1)[1].strip()
                    try:
                        return conv(text)
                    except ValueError:
                        raise ValueError(f"{path}:{n}: {section}.{key} '{text}' (expected "
                                         f"{'an integer' if conv is int else 'a number'})")
    except OSError:
        pass
    return default
