"""What the study plots share: matplotlib's pyplot, or a note without it."""


def pyplot_or_note(source):
    """pyplot with the file backend, or None after printing why no plot is
    written (the numbers stay in `source`)."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("note: matplotlib is not installed (apt-get install python3-matplotlib); no plot written,"
              f" the numbers are in {source}")
        return None
    return plt
