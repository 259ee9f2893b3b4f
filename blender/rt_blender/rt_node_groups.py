"""Shader nodes inside node groups, seen as Blender evaluates them: a node inside a group is
a `GroupNode` that remembers the group nodes it was reached through, and its sockets'
links and values are those of the tree around the group where they come from its Group
Input (a value the group node's socket holds, or whatever is linked into it there), and
those of the nodes inside where they come from another group's output. Reroutes are
passed through and muted links not followed, as Blender evaluates them; muted nodes are
left to the code that reads the links.

rt_shader_nodes, rt_shader_graphs and rt_export read a `GroupNode` as they read a node
(`type`, `inputs["Base Color"]`, `default_value`, `links[0].from_node`, …): the export
follows a material's surface into a group (a Principled BSDF in an asset's group, a Mix of
shaders a group makes) with no change to what it does outside one. Only baking, which
edits the material's own tree, stops at a group (warned).
"""


def _output_index(node, socket):
    return next(i for i, s in enumerate(node.outputs) if s == socket)


def active_output(tree, kind="GROUP_OUTPUT"):
    """A tree's active output node of type `kind` (its first if none is marked), or None."""
    outputs = [n for n in tree.nodes if n.type == kind]
    return next((n for n in outputs if getattr(n, "is_active_output", False)), outputs[0] if outputs else None)


class Link:
    """A link as seen from inside the groups: `from_node` and `from_socket` wrapped."""

    is_muted = False

    def __init__(self, from_socket, groups, to_socket):
        self.from_node = wrap_node(from_socket.node, groups)
        self.from_socket = GroupSocket(from_socket, groups, self.from_node)
        self.to_socket = to_socket


def resolve(socket, groups):
    """What feeds input `socket` (inside `groups`, outermost first): ("link", Link) or
    ("value", the value of the socket that holds it)."""
    links = [link for link in socket.links if not link.is_muted]
    if not links:
        return "value", socket
    link = links[0]
    node = link.from_node
    if node.type == "REROUTE":
        return resolve(node.inputs[0], groups)
    if node.type == "GROUP_INPUT" and groups:
        outer = groups[-1].inputs[_output_index(node, link.from_socket)]
        return resolve(outer, groups[:-1])
    if node.type == "GROUP" and node.node_tree is not None:
        inner = active_output(node.node_tree)
        if inner is None:
            return "value", None
        return resolve(inner.inputs[_output_index(node, link.from_socket)], groups + (node,))
    return "link", Link(link.from_socket, groups, socket)


class GroupSocket:
    """A socket of a node reached through `groups`: its links and value resolved."""

    def __init__(self, socket, groups, node):
        self.socket, self.groups, self.node = socket, groups, node

    def __getattr__(self, name):
        return getattr(self.socket, name)

    def __eq__(self, other):
        return isinstance(other, GroupSocket) and (self.socket, self.groups) == (other.socket, other.groups)

    def __hash__(self):
        return hash((self.socket.as_pointer(), tuple(g.as_pointer() for g in self.groups)))

    def _source(self):
        if self.socket.is_output:
            return "value", self.socket
        return resolve(self.socket, self.groups)

    @property
    def links(self):
        kind, what = self._source()
        return [what] if kind == "link" else []

    @property
    def is_linked(self):
        return self._source()[0] == "link"

    @property
    def default_value(self):
        kind, what = self._source()
        if kind == "value" and what is not None and hasattr(what, "default_value"):
            return what.default_value
        return self.socket.default_value


class Sockets:
    """A node's inputs or outputs, wrapped: by name, by place, `get`, `in`, iteration."""

    def __init__(self, sockets, node):
        self.sockets, self.node = sockets, node

    def _wrap(self, socket):
        return GroupSocket(socket, self.node.groups, self.node)

    def __getitem__(self, key):
        return self._wrap(self.sockets[key])

    def get(self, key, default=None):
        socket = self.sockets.get(key)
        return default if socket is None else self._wrap(socket)

    def __contains__(self, key):
        return key in self.sockets

    def __iter__(self):
        return (self._wrap(s) for s in self.sockets)

    def __len__(self):
        return len(self.sockets)


class GroupNode:
    """A node reached through the group nodes `groups` (outermost first)."""

    def __init__(self, node, groups):
        self.node, self.groups = node, groups
        self.inputs, self.outputs = Sockets(node.inputs, self), Sockets(node.outputs, self)

    def __getattr__(self, name):
        return getattr(self.node, name)

    def __eq__(self, other):
        return isinstance(other, GroupNode) and (self.node, self.groups) == (other.node, other.groups)

    def __hash__(self):
        return hash((self.node.as_pointer(), tuple(g.as_pointer() for g in self.groups)))


def wrap_node(node, groups):
    """`node` as reached through `groups`: itself outside any group."""
    return GroupNode(node, groups) if groups else node


def linked_node(socket):
    """The node linked into input `socket`, through node groups (entering a group whose
    output it is, leaving one through its Group Input), or None."""
    if isinstance(socket, GroupSocket):
        links = socket.links
        return links[0].from_node if links else None
    kind, what = resolve(socket, ())
    return what.from_node if kind == "link" else None


def followed(socket):
    """Input `socket` with its links followed through node groups (itself if it already is)."""
    if isinstance(socket, GroupSocket):
        return socket
    return GroupSocket(socket, (), socket.node)


def unwrap(socket, groups=()):
    """(the socket, the group nodes around it) for code that walks groups itself."""
    if isinstance(socket, GroupSocket):
        return socket.socket, socket.groups + tuple(groups)
    return socket, groups


def in_group(thing):
    """Whether a node or socket was reached inside a node group."""
    return bool(getattr(thing, "groups", ()))
