"""springnet"""
