angle factor: 8
function: cpfg_vocabulary.func 100
