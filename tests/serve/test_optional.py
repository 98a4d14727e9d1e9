from homesim.serve import optional


def test_missing_module_is_reported_not_raised():
    function, why = optional._optional_function("homesim.no_such_module", "f")
    assert function is None and "homesim.no_such_module is not available" in why


def test_missing_function_is_reported():
    function, why = optional._optional_function("homesim.program", "no_such_function")
    assert function is None and why == "homesim.program has no no_such_function()"


def test_present_function_is_returned():
    function, why = optional._optional_function("homesim.program", "parse_program")
    assert callable(function) and why == ""
