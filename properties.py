"""scene.fibrilfit: the sidebar's parameters, made from the one parameter definition."""
CLASSES = ()


def attach():
    pass


def detach():
    pass
