angle increment: 20
