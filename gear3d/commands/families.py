"""``gear3d families``: list the profile families."""


def add_parser(sub):
    return sub.add_parser("families", help="list gear families")


def run(args) -> int:
    from ..profiles import families
    print("\n".join(families()))
    return 0
