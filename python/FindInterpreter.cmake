# Which python3 the package is built for and tested with. The Debian packages it is used with
# (python3-numpy, -pandas, -matplotlib, -pytest) belong to one interpreter; a python3 earlier on
# PATH (pyenv, a virtual environment) may lack them, and testing there would skip what CI must run.
# So the first of "python3 on PATH, /usr/bin/python3" that imports numpy and pytest is chosen;
# -DPython_EXECUTABLE=... overrides.
if(NOT Python_EXECUTABLE)
  find_program(CHUTELAB_PATH_PYTHON3 python3)
  set(_chutelab_python "")
  foreach(candidate IN ITEMS ${CHUTELAB_PATH_PYTHON3} /usr/bin/python3)
    if(EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import numpy, pytest"
                      RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
      if(rc EQUAL 0)
        set(_chutelab_python "${candidate}")
        break()
      endif()
    endif()
  endforeach()
  if(NOT _chutelab_python AND CHUTELAB_PATH_PYTHON3)
    set(_chutelab_python "${CHUTELAB_PATH_PYTHON3}")
  endif()
  if(_chutelab_python)
    set(Python_EXECUTABLE "${_chutelab_python}" CACHE FILEPATH "python3 the package is built for")
  endif()
endif()
# pybind11 then finds that interpreter's headers through CMake's FindPython.
set(PYBIND11_FINDPYTHON ON)
