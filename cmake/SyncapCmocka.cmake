# syncap_cmocka_test(<name> LABEL unit|hil SOURCES ... [LIBS ...]) is defined here (firmware tests).
